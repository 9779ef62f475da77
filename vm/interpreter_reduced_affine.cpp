// vm/interpreter_reduced_affine.cpp: Interpreter<ReducedAffine>, instantiated from the one loop in interpreter.inl.
#include "vm/interpreter.inl"

namespace affray::vm {
template class Interpreter<ReducedAffine>;
}  // namespace affray::vm
