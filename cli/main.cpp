#include "cli/app.h"
#include "cli/heap_tuning.h"

int main(int argc, char** argv) {
  lcs::tune_heap_for_simulation();
  return lcs::run_cli(argc, argv);
}
