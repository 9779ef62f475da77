// vm/interpreter_affine.cpp: Interpreter<Affine>, instantiated from the one loop in interpreter.inl.
#include "vm/interpreter.inl"

namespace affray::vm {
template class Interpreter<Affine>;
}  // namespace affray::vm
