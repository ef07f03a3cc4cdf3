"""Scene files (TOML) shipped with upliftlab: the cases of Ewing's study and more."""
