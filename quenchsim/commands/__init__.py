"""Handlers of the top-level CLI commands (argument parsing + calls into the library)."""
