"""Reporting: text reports and plots of finished results (never a model run)."""
