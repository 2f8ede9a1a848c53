"""biceps: a shaded 3D biceps in the terminal, at exactly constant volume.

One namespace for three parts: ``biceps.engine`` (the model and the picture, no terminal),
``biceps.tui`` (the Textual app) and ``biceps.configs`` (the bundled models), with the
command line, ``biceps.cli``, above both.
"""
