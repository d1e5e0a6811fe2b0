# bench/local.mk: benchmark tooling. gen_scene writes scenes of a given
# triangle count, cavalry_bench measures load/BVH/render with GL timer
# queries, plot draws convergence curves; `make bench` runs bench/run.sh.
noinst_PROGRAMS += bench/gen_scene bench/plot
bench_gen_scene_SOURCES = bench/gen_scene.c
bench_gen_scene_LDADD = -lm
bench_plot_SOURCES = bench/plot.c
bench_plot_LDADD = $(PNG_LIBS) $(ZLIB_LIBS) -lm
noinst_PROGRAMS += bench/cavalry_bench
bench_cavalry_bench_SOURCES = bench/cavalry_bench.c bench/bench.h bench/record.c \
	bench/stages.c bench/summarize.c
bench_cavalry_bench_LDADD = $(CV_LIBS)
bench_cavalry_bench_CPPFLAGS = $(AM_CPPFLAGS) -I$(top_srcdir)/glsl
# veach-mis: direct light on the plates, computed independently of the GLSL
noinst_PROGRAMS += bench/mis_direct
bench_mis_direct_SOURCES = bench/mis_direct.c
bench_mis_direct_LDADD = $(CV_LIBS) -lm

# `make bench`: the quick set (minutes on llvmpipe) against this build tree.
# Full sizes, e.g. on the GPU machine: bench/run.sh --binary bench/cavalry_bench
.PHONY: bench
bench: bench/cavalry_bench bench/gen_scene
	$(SHELL) $(srcdir)/bench/run.sh --quick --binary bench/cavalry_bench \
		--work bench/out --out bench/out/quick.json

EXTRA_DIST += bench/common.sh bench/run.sh bench/converge.sh bench/csv_median.sh bench/coldstart.sh \
	bench/guiding.sh bench/README.md \
	bench/RESULTS.md
TESTS += bench/bench_test.sh
EXTRA_DIST += bench/bench_test.sh

# `make bench-multigpu`: the wall time of N jobs on GPU 0, then on every GPU
# (bench/multigpu.sh; its options through MULTIGPU_FLAGS, e.g. "--jobs 32").
.PHONY: bench-multigpu
bench-multigpu: src/cavalry-batch bench/gen_scene
	$(SHELL) $(srcdir)/bench/multigpu.sh --binary src/cavalry-batch $(MULTIGPU_FLAGS)
EXTRA_DIST += bench/multigpu.sh bench/bdpt.sh
# the register proxy of shade kernels (bench/amd_regs/stats.sh: RADV, no GPU)
EXTRA_DIST += bench/amd_regs/stats.sh bench/amd_regs/assemble.c bench/amd_regs/vkstats.c bench/amd_regs/remap.py
# the CPU time of rlpath sdtree's host refinement from splatted statistics
noinst_PROGRAMS += bench/sdtree_build
bench_sdtree_build_SOURCES = bench/sdtree_build.c
bench_sdtree_build_LDADD = $(CV_LIBS) -lm
# traversal work per ray (nodes, triangles) of the GPU-built tree on a scene
noinst_PROGRAMS += bench/bvh_work
bench_bvh_work_SOURCES = bench/bvh_work.c bench/rays.c bench/rays.h bench/scene_tree.c \
	bench/scene_tree.h tests/bvh/sah_ref.h tests/bvh/widen_ref.h
bench_bvh_work_LDADD = $(CV_LIBS) -lm
bench_bvh_work_CPPFLAGS = $(AM_CPPFLAGS) -I$(top_srcdir)/glsl
# the same rays on Cavalry's traversal and on the RT cores (Vulkan
# ray-tracing pipelines); built only where configure found Vulkan and
# glslangValidator. The shaders' SPIR-V is compiled into the binary.
RT_PROBE_SPV = bench/rt_probe_rgen.h bench/rt_probe_rchit.h bench/rt_probe_rmiss.h
EXTRA_DIST += bench/rt_probe.rgen bench/rt_probe.rchit bench/rt_probe.rmiss \
	bench/rt_probe_payload.glsl
if HAVE_RT_PROBE
noinst_PROGRAMS += bench/rt_probe
bench_rt_probe_SOURCES = bench/rt_probe.c bench/rays.c bench/rays.h bench/scene_tree.c \
	bench/scene_tree.h bench/rt_vk.c bench/rt_vk.h
nodist_bench_rt_probe_SOURCES = $(RT_PROBE_SPV)
bench_rt_probe_LDADD = $(CV_LIBS) $(VULKAN_LIBS) -lm
bench_rt_probe_CPPFLAGS = $(AM_CPPFLAGS) -I$(top_srcdir)/glsl $(VULKAN_CFLAGS)
BUILT_SOURCES += $(RT_PROBE_SPV)
bench/rt_probe-rt_vk.$(OBJEXT): $(RT_PROBE_SPV)
CLEANFILES += $(RT_PROBE_SPV)
# bench/rt_probe.STAGE -> bench/rt_probe_STAGE.h: a uint32_t array named
# rt_probe_STAGE (glslangValidator prints its messages on stdout: shown
# only when it fails)
bench/rt_probe_%.h: $(srcdir)/bench/rt_probe.% $(srcdir)/bench/rt_probe_payload.glsl
	@$(MKDIR_P) bench
	$(AM_V_GEN)$(GLSLANG) --target-env vulkan1.2 -V --vn rt_probe_$* -o $@.tmp $< >$@.log 2>&1 \
		|| { cat $@.log; rm -f $@.log $@.tmp; exit 1; }; rm -f $@.log; mv $@.tmp $@
endif
