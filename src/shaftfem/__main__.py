from shaftfem.cli import entry

entry()
