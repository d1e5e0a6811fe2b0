# contrib/: files for farm schedulers, installed with the documentation for
# people to copy and adapt (tests/contrib checks them).
slurmdocdir = $(docdir)/slurm
dist_slurmdoc_DATA = contrib/slurm/README.md contrib/slurm/cavalry.sbatch
k8sdocdir = $(docdir)/k8s
dist_k8sdoc_DATA = contrib/k8s/README.md contrib/k8s/cavalry-job.yaml
