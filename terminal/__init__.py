"""The terminal layer: what the terminal can show, and pictures written in its protocols,
free of Textual (the app and ``biceps snapshot`` alike use it)."""
