# src/output: see Makefile.am
