# src/manifest: see Makefile.am
