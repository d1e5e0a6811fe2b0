# src/bvh: GPU BVH build (LBVH + treelet restructuring) and traversal GLSL.
libcavalry_a_SOURCES += \
	src/bvh/bounds.c src/bvh/bounds.h \
	src/bvh/bvh.c src/bvh/bvh.h src/bvh/curve_bvh.c src/bvh/curve_bvh.h \
	src/bvh/median_split.c src/bvh/median_split.h \
	src/bvh/motion_bvh.c src/bvh/motion_bvh.h \
	src/bvh/radix_sort.c src/bvh/radix_sort.h \
	src/bvh/scan.c src/bvh/scan.h \
	src/bvh/scratch.c src/bvh/scratch.h \
	src/bvh/split.c src/bvh/split.h \
	src/bvh/treelet_schedule.c src/bvh/treelet_schedule.h \
	src/bvh/widen.c src/bvh/widen.h

GLSL_FILES += \
	glsl/shared/bvh.h \
	glsl/bvh/bounds.comp glsl/bvh/morton.comp \
	glsl/bvh/radix_digits.glsl glsl/bvh/radix_count.comp glsl/bvh/radix_spine.comp \
	glsl/bvh/radix_scatter.comp \
	glsl/bvh/scan_block.comp glsl/bvh/scan_add.comp \
	glsl/bvh/hierarchy.comp glsl/bvh/refit.comp glsl/bvh/sah.glsl glsl/bvh/treelet.comp \
	glsl/bvh/layout.comp glsl/bvh/emit.comp glsl/bvh/leaf_tris.comp glsl/bvh/leaf_slots.comp \
	glsl/bvh/split.glsl glsl/bvh/split_priority.comp \
	glsl/bvh/split_sum.comp glsl/bvh/split_count.comp glsl/bvh/split_emit.comp \
	glsl/bvh/split_remap.comp \
	glsl/bvh/widen.glsl glsl/bvh/widen_next.comp glsl/bvh/widen_level.comp \
	glsl/bvh/widen_emit.comp glsl/bvh/widen_up.comp glsl/bvh/widen_cost.comp \
	glsl/bvh/mesh_buffers.glsl glsl/bvh/scene_buffers.glsl glsl/bvh/triangle.glsl glsl/bvh/traverse.glsl \
	glsl/bvh/rays_test.comp glsl/bvh/curves_test.comp \
	glsl/bvh/motion.glsl glsl/bvh/motion_test.comp
