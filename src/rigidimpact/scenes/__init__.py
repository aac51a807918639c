"""The scene format (TOML) and its one reader."""
