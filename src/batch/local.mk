# src/batch: see Makefile.am
