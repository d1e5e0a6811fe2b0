# src/scene: see Makefile.am
