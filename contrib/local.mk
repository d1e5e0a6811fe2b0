# contrib/: files for farm schedulers, installed with the documentation for
# people to copy and adapt (tests/contrib checks them).
slurmdocdir = $(docdir)/slurm
dist_slurmdoc_DATA = contrib/slurm/README.md contrib/slurm/cavalry.sbatch
