"""The case and its physics: validated parameters, initial shapes and defects, the radiation load,
the closed-form theory of the paper's Section II and exact results for the discrete chain."""
