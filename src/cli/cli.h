/* cli.h: the command line of cavalry-batch (getopt_long); returns the
 * process exit status documented in cavalry-batch(1). */
#ifndef CV_CLI_CLI_H
#define CV_CLI_CLI_H

int cv_cli_main(int argc, char **argv);

#endif
