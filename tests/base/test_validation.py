"""The one-line error of a bad value (base.validation): the value as a user reads it, as the help writes it."""

import numpy as np
import pytest

from lightsail_mbs.base.validation import ParameterError, check, finite


@pytest.mark.parametrize(
    "value, text",
    [(1e9, "1e+09"), (-1e8, "-1e+08"), (np.float64(0.3), "0.3"), (2.5e-7, "2.5e-07"), (3, "3"), ("x", "'x'")],
)
def test_a_refused_value_is_written_as_a_user_reads_it(value, text):
    with pytest.raises(ParameterError) as err:
        check("field", value, False, "something else")
    assert str(err.value) == f"field={text} is invalid: allowed something else"


def test_a_value_that_is_not_finite_is_named_in_one_line():
    with pytest.raises(ParameterError, match=r"^field=inf is invalid: allowed a finite real number \(no NaN or inf\)$"):
        finite("field", float("inf"))
    with pytest.raises(ParameterError, match="^field='1' is invalid: allowed a finite real number$"):
        finite("field", "1")
