# man/local.mk
dist_man_MANS += man/cavalry-manifest.5
