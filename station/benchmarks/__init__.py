"""Benchmarks behind ``station bench``; shared report writing in ``report.py``."""
