// vm/interpreter_dual_interval.cpp: Interpreter<Dual<Interval>>, for interval bounds of shaders
// that take derivatives. Instantiated from the one loop in interpreter.inl.
#include "vm/interpreter.inl"

namespace affray::vm {
template class Interpreter<Dual<Interval>>;
}  // namespace affray::vm
