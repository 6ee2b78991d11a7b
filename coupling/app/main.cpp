// The tmdem program: contract section 1. Everything is in tmdem_main (coupling/app/TmdemMain.h).
#include "coupling/app/TmdemMain.h"

int main(int argc, char** argv) { return tmdem::coupling::tmdem_main(argc, argv); }
