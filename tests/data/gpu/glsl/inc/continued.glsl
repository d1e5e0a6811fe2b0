// continued.glsl: a #define continued over lines in an included file.
#define PAIR_SUM \
    (4.0 + 5.0)
