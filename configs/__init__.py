"""The bundled models, installed as package data and read through ``importlib.resources``."""
