// vm/interpreter_dual.cpp: Interpreter<Dual<double>>, instantiated from the one loop in interpreter.inl.
#include "vm/interpreter.inl"

namespace affray::vm {
template class Interpreter<Dual<double>>;
}  // namespace affray::vm
