# tests/gpu: see tests/local.mk
