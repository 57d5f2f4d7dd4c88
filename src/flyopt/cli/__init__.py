"""The command line: one argparse tree and one exit-code table."""
