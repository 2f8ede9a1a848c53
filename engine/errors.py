"""The errors the engine raises on purpose, each carrying a message a person can act on."""


class BicepsError(Exception):
    """Base of every deliberate refusal: the message is meant for the user as it is."""


class RefusedChange(BicepsError):
    """A change to the model was refused; the model is left exactly as it was."""


class ConfigError(BicepsError):
    """A configuration file cannot be read, validated or written."""


class SettingError(BicepsError):
    """A view, light or render setting outside its rules: no such setting was made."""


class FileError(BicepsError):
    """A file cannot be read or written; whatever was there before is untouched."""


class FileChanged(FileError):
    """The file was changed on disk since it was read: saving would lose those changes."""


def shown(text: str) -> str:
    """What a person typed, as a message quotes it: ``'abc'``, or ``nothing``."""
    return repr(text.strip()) if text.strip() else "nothing"
