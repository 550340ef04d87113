#error "LCM in an algorithm library: algorithms take plain C++ types; only nodes (*_node.cc, *_main.cc) and tools may include LCM."
