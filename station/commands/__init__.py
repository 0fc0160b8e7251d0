"""One module per ``station`` subcommand; see ``station.cli``."""
