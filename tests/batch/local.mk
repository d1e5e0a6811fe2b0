# tests/batch: see tests/local.mk
