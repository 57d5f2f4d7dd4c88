"""Input: scene files (TOML, with units) to a Scene."""
