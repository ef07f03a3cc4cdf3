"""upliftlab.reduced"""
