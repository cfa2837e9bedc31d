// Translation unit for library folders that have no sources yet (keeps CMake targets valid).
