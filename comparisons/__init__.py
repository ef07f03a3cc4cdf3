"""upliftlab.comparisons"""
