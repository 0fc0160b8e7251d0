"""Camera and line I/O drivers. Imports without torch."""
