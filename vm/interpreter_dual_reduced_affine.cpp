// vm/interpreter_dual_reduced_affine.cpp: Interpreter<Dual<ReducedAffine>>, instantiated from the one loop in interpreter.inl.
#include "vm/interpreter.inl"

namespace affray::vm {
template class Interpreter<Dual<ReducedAffine>>;
}  // namespace affray::vm
