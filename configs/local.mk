# configs/: the OpenColorIO config Cavalry ships. It is also compiled into
# the binary (src/color/embed_config.sh); the installed copy is for people
# to read, copy and point color.config or $OCIO at.
configsdir = $(pkgdatadir)/configs
dist_configs_DATA = configs/cavalry.ocio
EXTRA_DIST += configs/example/manifest.yaml configs/example/scene.pbrt
