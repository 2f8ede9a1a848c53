"""The app's screens: the main one, help, and the dialogs."""
