"""The main screen's widgets: the picture, the node table and the numbers."""
