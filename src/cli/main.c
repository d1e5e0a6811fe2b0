/* main.c: entry point of cavalry-batch. Parses the command line and hands
 * the work to the batch stage; the only place that decides the exit status. */
#include "cli/cli.h"

int main(int argc, char **argv)
{
    return cv_cli_main(argc, argv);
}
