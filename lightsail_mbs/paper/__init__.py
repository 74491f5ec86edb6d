"""The pipelines behind the paper's figures, importable so that a regular install reproduces them."""
