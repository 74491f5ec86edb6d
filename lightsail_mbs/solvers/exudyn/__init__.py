"""The Exudyn solver: the chain as one ObjectKinematicTree integrated by Exudyn."""
