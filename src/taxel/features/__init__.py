"""Passive tactile features of one tactile image (Ellis seed, section 2.1)."""
