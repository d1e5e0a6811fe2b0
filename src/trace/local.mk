# src/trace: see Makefile.am
