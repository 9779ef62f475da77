// vm/interpreter_interval.cpp: Interpreter<Interval>, instantiated from the one loop in interpreter.inl.
#include "vm/interpreter.inl"

namespace affray::vm {
template class Interpreter<Interval>;
}  // namespace affray::vm
