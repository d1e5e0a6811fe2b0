# src/gpu: see Makefile.am
