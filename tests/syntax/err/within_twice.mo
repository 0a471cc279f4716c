within A;
within B;
model M
end M;
