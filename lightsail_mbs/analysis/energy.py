"""Energy of a run: kinetic plus elastic energy and the heat of the dampers (defined in
:mod:`lightsail_mbs.model.energy`, which the Result's summary uses; importable from here too)."""

from lightsail_mbs.model.energy import dissipated_energy, dissipated_power, mechanical_energy

__all__ = ["dissipated_energy", "dissipated_power", "mechanical_energy"]
