"""The terminal app around the engine: Textual screens, widgets and keys."""
