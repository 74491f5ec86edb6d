"""The case and its physics: validated parameters, initial shapes and defects, the radiation load and the
other physics terms every solver applies (:mod:`lightsail_mbs.model.terms`), the closed-form theory of the
paper's Section II and exact results for the discrete chain."""
