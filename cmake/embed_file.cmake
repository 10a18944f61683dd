# cmake -DIN=file.cl -DOUT=file.cpp -DSYMBOL=name -P embed_file.cmake
file(READ "${IN}" content HEX)
string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${content}")
file(WRITE "${OUT}.tmp"
  "// Generated from ${IN}; do not edit.\nnamespace isocurv { namespace kernels {\n"
  "static const char ${SYMBOL}_data[] = {${bytes} 0x00};\n"
  "extern const char* const ${SYMBOL};\nconst char* const ${SYMBOL} = ${SYMBOL}_data;\n} }\n")
file(RENAME "${OUT}.tmp" "${OUT}")
