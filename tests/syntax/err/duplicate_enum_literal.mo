type State = enumeration(Flight, Sliding, Flight);
