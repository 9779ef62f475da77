/* tests/tools/check_layers/lang/parser.y: the C++ blocks of a Bison source are checked too: lang/
   includes diag/, and a generated header beside it, but not texture/, which it does not link. */
%code requires {
#include "diag/diagnostic.h"
#include "lang/ast.h"
#include "texture/texture.h"  // crosses the layers
}
%{
#include "parser.hh"
%}
%%
unit: ;
%%
