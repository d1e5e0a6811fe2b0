# tests/trace: see tests/local.mk
