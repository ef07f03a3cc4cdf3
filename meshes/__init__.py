"""upliftlab.meshes"""
