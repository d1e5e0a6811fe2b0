// fine.glsl: compiles.
void fine() {}
