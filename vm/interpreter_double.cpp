// vm/interpreter_double.cpp: Interpreter<double>, instantiated from the one loop in interpreter.inl.
#include "vm/interpreter.inl"

namespace affray::vm {
template class Interpreter<double>;
}  // namespace affray::vm
