# A touch probe (di1) for search_di.mod: TIME SIGNAL VALUE, robot time in seconds.
3.0 di1 1
3.5 di1 0
6.0 di1 1
