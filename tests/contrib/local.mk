# tests/contrib: the farm scheduler files under contrib/ (Slurm, Kubernetes).
TESTS += tests/contrib/slurm_test.sh tests/contrib/k8s_test.sh
EXTRA_DIST += tests/contrib/slurm_test.sh tests/contrib/k8s_test.sh tests/contrib/k8s_check.py \
	tests/data/batch/five.yaml
