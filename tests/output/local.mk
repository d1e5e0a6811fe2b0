# tests/output: see tests/local.mk
