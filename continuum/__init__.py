"""upliftlab.continuum"""
