# tests/manifest: see tests/local.mk
