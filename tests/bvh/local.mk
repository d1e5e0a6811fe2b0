# tests/bvh: see tests/local.mk
