/* cli.c: placeholder until the gpu stage lands (replaced below). */
#include "cli/cli.h"
int cv_cli_main(int argc, char **argv) { (void)argc; (void)argv; return 0; }
