"""The in-house reduced-Lagrangian solver, independent of Exudyn."""
