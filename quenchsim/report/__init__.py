"""Plots and the Markdown/HTML reports (quench validation pages and bearing-module pages)."""
