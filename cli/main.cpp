#include "cli/app.h"

int main(int argc, char** argv) { return lcs::run_cli(argc, argv); }
