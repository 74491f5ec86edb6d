"""Pictures of Results: the scene of a frame, its two canvases (Exudyn's raytracer, matplotlib),
frames and movies, and the recurring plots on matplotlib's object API."""
