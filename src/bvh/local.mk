# src/bvh: see Makefile.am
