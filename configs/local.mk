# configs/local.mk
