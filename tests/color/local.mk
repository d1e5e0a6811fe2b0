# tests/color: see tests/local.mk
