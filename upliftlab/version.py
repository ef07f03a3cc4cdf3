"""upliftlab's version, apart so that any module can name it without importing the package's
face (which loads the numba cache settings)."""

__version__ = "0.1.0"
