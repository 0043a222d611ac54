"""Labelling: which dictionary object a region is (colour and shape, OpenCLIP), and the
VLM path that asks a vision-language model for the whole graph instead.
"""
