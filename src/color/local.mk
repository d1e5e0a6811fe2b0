# src/color: see Makefile.am
