// vm/interpreter_dual_affine.cpp: Interpreter<Dual<Affine>>, instantiated from the one loop in interpreter.inl.
#include "vm/interpreter.inl"

namespace affray::vm {
template class Interpreter<Dual<Affine>>;
}  // namespace affray::vm
